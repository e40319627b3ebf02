// models.h: the analytic layered models gonio compares with the reference, all of host/models but the comparison
// (compare.h): the registry (model_registry.h), which stacks each represents (model_applicability.h), their bin
// averages on the device (model_evaluator.h) and how each term is integrated (model_plan.h), the CPU twin
// (model_cpu.h), Belcour's tables (belcour_tables_host.h) and the models' per-stack tables (stack_tables.h).
#pragma once
#include "belcour_tables_host.h"
#include "stack_tables.h"
#include "model_applicability.h"
#include "model_cpu.h"
#include "model_evaluator.h"
#include "model_plan.h"
#include "model_registry.h"

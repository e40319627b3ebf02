// cmd_models.h: `gonio models`: the models' ids, citations, and which stacks each represents.
#pragma once

namespace gonio {

int cmd_models();

}   // namespace gonio

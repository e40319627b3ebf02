// python_tool.h: the figures and HTML pages, drawn by gonio's Python tools (tools/*.py).
#pragma once
#include <string>
#include <vector>

namespace gonio {

// Runs tools/<script> DIR with python_interpreter();
// warns (naming `what`) if it fails: the numbers are written already. Compare's report, bench's and sweep's figures.
void run_python_tool(const std::string& script, const std::string& dir, const std::string& what);

// Runs tools/<script> ARGS... with the same Python and returns its exit status (127 if it could not start).
int run_python_command(const std::string& script, const std::vector<std::string>& args);

// The Python that runs the tools: GONIO_PYTHON, else the venv beside the gonio binary (./run test makes it, with
// OpenEXR and mitsuba), else /usr/bin/python3, else python3 on the PATH.
std::string python_interpreter();

}   // namespace gonio

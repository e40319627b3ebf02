// python_tool.h: the figures and HTML pages, drawn by gonio's Python tools (tools/*.py).
#pragma once
#include <string>

namespace gonio {

// Runs tools/<script> DIR with Python 3 (GONIO_PYTHON, else /usr/bin/python3, else python3 on the PATH);
// warns (naming `what`) if it fails: the numbers are written already. Compare's report, bench's and sweep's figures.
void run_python_tool(const std::string& script, const std::string& dir, const std::string& what);

}  // namespace gonio

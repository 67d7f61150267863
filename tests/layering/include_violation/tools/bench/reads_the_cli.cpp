// Fixture of tests/layering/layering_checks.sh: a benchmark engine that includes the command line.
#include "tools/cli/commands.hpp"

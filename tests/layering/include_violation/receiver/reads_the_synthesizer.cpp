// Fixture of tests/layering/layering_checks.sh: a receiver source that includes the synthesizer.
#include "signals/sim/if_synthesizer.hpp"

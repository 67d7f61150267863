"""Assertions of single command-line tests (tests/cli/NAME.sh runs checks.NAME), each a
list of named checks over that test's products."""

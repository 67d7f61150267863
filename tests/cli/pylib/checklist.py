"""Named checks of one test step: each prints ok or FAIL with the value it judged, and the
step exits non-zero when any failed."""
import sys


class CheckList:
    def __init__(self, prefix=""):
        self.prefix = prefix + ": " if prefix else ""
        self.failed = 0

    def check(self, name, ok, value=""):
        print(("ok   " if ok else "FAIL ") + self.prefix + name, value)
        self.failed += not ok
        return ok

    def exit(self):
        sys.exit(1 if self.failed else 0)

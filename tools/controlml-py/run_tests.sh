#!/usr/bin/env bash
# Runs controlml.py's unit tests (codec against docs/CONTROLML.md's examples, slixmpp wire form, arguments) in its
# venv (created on first use by venv.sh). Last line: "controlml-py: N passed, N failed". Exit 0 only when all pass.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
python=$("$here/venv.sh")
cd "$here"
exec "$python" - <<'PY'
import sys, unittest
result = unittest.TextTestRunner(verbosity=1).run(unittest.defaultTestLoader.discover("tests"))
failed = len(result.failures) + len(result.errors) + len(result.unexpectedSuccesses)
skipped = len(result.skipped)
print(f"controlml-py: {result.testsRun - failed - skipped} passed, {failed + skipped} failed")
sys.exit(0 if failed == 0 and skipped == 0 and result.testsRun > 0 else 1)
PY

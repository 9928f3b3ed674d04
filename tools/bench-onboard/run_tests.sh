#!/usr/bin/env bash
# Runs bench_onboard.py's unit tests (its report against log lines formatted from the onboard's Java sources) in
# controlml.py's venv. Last line: "bench-onboard: N passed, N failed". Exit 0 only when all pass.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
python=$("$here/../controlml-py/venv.sh")
cd "$here"
exec "$python" - <<'PY'
import sys, unittest
result = unittest.TextTestRunner(verbosity=1).run(unittest.defaultTestLoader.discover("tests"))
failed = len(result.failures) + len(result.errors) + len(result.unexpectedSuccesses)
skipped = len(result.skipped)
print(f"bench-onboard: {result.testsRun - failed - skipped} passed, {failed + skipped} failed")
sys.exit(0 if failed == 0 and skipped == 0 and result.testsRun > 0 else 1)
PY

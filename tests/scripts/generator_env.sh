# Sourced by the tests that draw worlds with scripts/random_scenarios.py: sets `python`
# (Debian's, which has NumPy when python3-numpy is installed) and a temporary folder `out`
# removed on exit; exits 77 (skipped) without NumPy.
python=/usr/bin/python3
"$python" -c "import numpy" 2>/dev/null || { echo "skipped: $python has no numpy (apt-get install python3-numpy)"; exit 77; }
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT

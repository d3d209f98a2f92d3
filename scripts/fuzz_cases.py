"""Runs fuzz cases, each in its own Python process with a time limit, so that a crash or a hang
is seen as such (the fuzz_*.py scripts share it)."""
import argparse
import subprocess
import sys
import time


def run_seeds(case_code, seeds, case_args, label, timeout):
    """Runs `case_code` (a Python program) for each seed with `case_args(seed)` as its arguments;
    prints one line per seed (`label(seed)`, then the case's last line of output, its exit or its
    time-out) and the failing seeds. Returns the process exit code: 1 if any seed failed."""
    failing = []
    for seed in seeds:
        t = time.perf_counter()
        try:
            p = subprocess.run([sys.executable, "-c", case_code, *map(str, case_args(seed))], capture_output=True,
                               text=True, timeout=timeout)
            if p.returncode != 0:
                failing.append(seed)
                last = (p.stdout.strip().splitlines() or p.stderr.strip().splitlines() or [""])[-1]
                status = f"FAILED (exit {p.returncode}): {last[:300]}"
            else:
                status = p.stdout.strip().splitlines()[-1][:300]
        except subprocess.TimeoutExpired as e:
            failing.append(seed)
            out = e.stdout.decode() if isinstance(e.stdout, bytes) else (e.stdout or "")
            status = f"TIMED OUT after {timeout:.0f} s: {(out.strip().splitlines() or [''])[-1][:300]}"
        print(f"seed {seed} ({label(seed)}): {status} [{time.perf_counter() - t:.1f} s]", flush=True)
    print("failing seeds:", failing or "none")
    return 1 if failing else 0


def seed_range(doc, timeout):
    """FIRST LAST [--timeout S] from the command line (`doc`: the script's docstring)."""
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    ap.add_argument("first", type=int)
    ap.add_argument("last", type=int, help="first seed not run (the range leaves it out)")
    ap.add_argument("--timeout", type=float, default=timeout)
    args = ap.parse_args()
    return range(args.first, args.last), args.timeout

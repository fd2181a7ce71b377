"""python3 -S -m exactinv_check CERT.json [CERT.json ...]

Exit status: 0 every certificate verified; 1 a claim was rejected (the last line says why: over the
kernel's budget, or a fault inside the kernel -- a bug, never an accept); 2 bad input (a file that
cannot be read or is not an exactinv certificate).  The kernel's own test: python3 -S -m exactinv_check.selftest."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from .kernel import check


def main(argv: Any = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python3 -S -m exactinv_check",
        description="The trusted kernel of exactinv: re-prove every claim of a certificate in exact "
                    "arithmetic, with the Python standard library only.",
        epilog="exit status: 0 verified, 1 rejected, 2 bad input")
    parser.add_argument("certificates", nargs="+", metavar="CERT.json")
    parser.add_argument("-q", "--quiet", action="store_true", help="print only the final verdict per file")
    args = parser.parse_args(argv)
    status = 0
    def progress(k: int, total: int, kind: str) -> None:
        if sys.stderr.isatty():
            print(f"\r  checking claim {k + 1}/{total}: {kind:<32}", end="", file=sys.stderr, flush=True)

    for path in args.certificates:
        report = check(path, progress)
        if sys.stderr.isatty():
            print("\r" + " " * 60 + "\r", end="", file=sys.stderr)
        text = str(report).splitlines()
        print(f"{path}:")
        print("\n".join(text[-1:] if args.quiet else text))
        status = max(status, 2 if report.bad_input else (0 if report.ok else 1))
    return status


if __name__ == "__main__":
    sys.exit(main())

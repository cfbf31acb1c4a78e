#!/usr/bin/env python3
"""Fails when a binary holds an AVX instruction (VEX/EVEX-encoded, or on ymm/zmm/mask registers:
AVX, AVX2, AVX-512) outside the functions allowed to (the dispatched kernels' AVX2 copies,
pss/KernelDispatch.cxx), so that the default build loads and runs on any x86-64 CPU (the baseline: SSE2).

    check_instructions.py [--objdump objdump] [--allow REGEX] [--kernels FILE]... [--v3 FILE]... FILE...

FILE may be an executable, a shared library or a static archive. A file given with --kernels is
checked too, and must also hold the allowed functions' AVX instructions (the dispatched copies
must exist where the core is linked in). A file given with --v3 (the core's copy for x86-64-v3)
is not checked for AVX; it must hold fused multiply-adds (vfmadd...), the proof that it was
compiled for x86-64-v3. Exit 0 when every file passes.
"""
import argparse
import re
import subprocess
import sys

FUNCTION = re.compile(r"^[0-9a-f]+ <(.+)>:$")
INSTRUCTION = re.compile(r"^\s+[0-9a-f]+:\s+(\S+)\s*(.*)$")
WIDE_REGISTER = re.compile(r"%(?:ymm|zmm)\d+|%k[0-7]\b")
NOT_AVX = {"verr", "verw"}


def avx_instructions(objdump, path):
    """Yields (function, instruction) for every AVX instruction in path."""
    out = subprocess.run([objdump, "-d", "-C", "--no-show-raw-insn", path], check=True,
                         stdout=subprocess.PIPE, universal_newlines=True).stdout
    function = "?"
    for line in out.splitlines():
        m = FUNCTION.match(line)
        if m:
            function = m.group(1)
            continue
        m = INSTRUCTION.match(line)
        if not m:
            continue
        mnemonic, operands = m.group(1), m.group(2)
        if (mnemonic.startswith("v") and mnemonic not in NOT_AVX) or WIDE_REGISTER.search(operands):
            yield function, (mnemonic + " " + operands).strip()


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--objdump", default="objdump")
    parser.add_argument("--allow", default=r"Avx2\b", help="regular expression on (demangled) function names")
    parser.add_argument("--kernels", action="append", default=[], help="a file that must hold the AVX2 copies")
    parser.add_argument("--v3", action="append", default=[], help="the core's copy for x86-64-v3")
    parser.add_argument("files", nargs="*")
    args = parser.parse_args()
    allow = re.compile(args.allow)
    failed = False
    for path in args.v3:
        fused = sum(1 for _, instruction in avx_instructions(args.objdump, path) if instruction.startswith("vfm"))
        if fused:
            print("ok   %s: %d fused multiply-adds (x86-64-v3)" % (path, fused))
        else:
            failed = True
            print("FAIL %s: no fused multiply-add: not compiled for x86-64-v3" % path)
    for path in args.kernels + args.files:
        offenders = {}
        allowed = set()
        for function, instruction in avx_instructions(args.objdump, path):
            if allow.search(function):
                allowed.add(function)
            else:
                offenders.setdefault(function, instruction)
        if offenders:
            failed = True
            print("FAIL %s: AVX instructions in %d function(s) outside the dispatched kernels:" % (path, len(offenders)))
            for function, instruction in sorted(offenders.items())[:20]:
                print("  %s: %s" % (function, instruction))
        elif path in args.kernels and not allowed:
            failed = True
            print("FAIL %s: no dispatched AVX2 kernel found (allowed: %s)" % (path, args.allow))
        else:
            print("ok   %s: baseline x86-64 outside %d dispatched function(s)" % (path, len(allowed)))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

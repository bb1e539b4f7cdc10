#!/usr/bin/env python3
"""Which objects of a static library a user of another static library pulls in when linking.

    check_link_closure.py [--nm NM] USER.a PROVIDER.a (--forbid NAME | --require NAME)...

Follows the undefined symbols of every object in USER.a through PROVIDER.a (as the linker does with archives:
an object is pulled when it defines a symbol still needed, and its own undefined symbols are needed in turn)
and checks the result: --forbid NAME fails when a pulled object defines a function whose demangled name starts
with NAME, --require NAME fails when none does. Exit code 0 when every check holds, 1 otherwise, 2 for bad use.
Used by CTest to show that rockfit::io does not link core's simulator while rockfit::synth does (docs/design.md §1).
"""
import argparse
import collections
import subprocess
import sys


def read_archive(path, nm):
    """member → (defined symbols, undefined symbols, demangled defined names), from `nm -A`."""
    members = collections.defaultdict(lambda: (set(), set(), set()))
    for demangle in (False, True):
        out = subprocess.run([nm, "-A"] + (["-C"] if demangle else []) + [path], capture_output=True, text=True,
                             check=True).stdout
        for line in out.splitlines():
            # "lib.a:member.o:ADDRESS T symbol" or "lib.a:member.o:          U symbol" (a symbol may hold spaces)
            head, _, rest = line.partition(" ")
            parts = head.split(":")
            fields = rest.strip().split(None, 1)
            if len(parts) < 3 or len(fields) != 2:
                continue
            member = parts[1]
            kind, symbol = fields
            if demangle:
                if kind in "TW":
                    members[member][2].add(symbol)
            elif kind == "U":
                members[member][1].add(symbol)
            elif kind in "TWDBRVui":
                members[member][0].add(symbol)
    return members


def pulled_objects(user, provider):
    defined_in = {}
    for member, (defined, _, _) in provider.items():
        for symbol in defined:
            defined_in.setdefault(symbol, member)
    own = set().union(*(d for d, _, _ in user.values())) if user else set()
    needed = [s for _, (_, undefined, _) in user.items() for s in undefined if s not in own]
    pulled, seen = set(), set()
    while needed:
        symbol = needed.pop()
        if symbol in seen:
            continue
        seen.add(symbol)
        member = defined_in.get(symbol)
        if member is not None and member not in pulled:
            pulled.add(member)
            needed.extend(provider[member][1])
    return pulled


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nm", default="nm", help="the nm program (default: nm from PATH)")
    parser.add_argument("user")
    parser.add_argument("provider")
    parser.add_argument("--forbid", action="append", default=[])
    parser.add_argument("--require", action="append", default=[])
    args = parser.parse_args()
    if not args.forbid and not args.require:
        parser.error("give at least one --forbid or --require")
    provider = read_archive(args.provider, args.nm)
    pulled = sorted(pulled_objects(read_archive(args.user, args.nm), provider))
    print(f"{args.user} pulls {len(pulled)} objects of {args.provider}: {' '.join(pulled) or 'none'}")
    def defines(name):
        return [m for m in pulled if any(f.startswith(name) for f in provider[m][2])]
    ok = True
    for name in args.forbid:
        where = defines(name)
        if where:
            print(f"FAIL: {name} is linked (defined in {' '.join(where)})")
            ok = False
    for name in args.require:
        if not defines(name):
            print(f"FAIL: {name} is not linked")
            ok = False
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())

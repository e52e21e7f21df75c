"""Rewrite tests/data/example_numbers.json: ``python -m tests.regenerate_example_numbers``
(from the repository root; a few minutes when the modal-data cache is cold).

Run it after a change that moves an example's numbers ON PURPOSE (a model change, an edited
example file), review the diff of the JSON file and commit it with the change. ``--only NAME``
(repeatable) recomputes the named cases and keeps the others.
"""

from __future__ import annotations

import argparse
import json

from .example_numbers import DATA, cases, compute, load_numbers


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", action="append", default=[], metavar="NAME",
                        help="a case to recompute (default: all)")
    args = parser.parse_args(argv)
    names = list(cases())
    unknown = sorted(set(args.only) - set(names))
    if unknown:
        parser.error(f"unknown cases {unknown}; known: {names}")
    numbers = load_numbers() if args.only else {}
    for name in args.only or names:
        numbers[name] = compute(name)
        print(f"{name}: {numbers[name]!r}", flush=True)
    ordered = {name: numbers[name] for name in names if name in numbers}
    DATA.parent.mkdir(parents=True, exist_ok=True)
    DATA.write_text(json.dumps(ordered, indent=2) + "\n")
    print(f"wrote {DATA}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

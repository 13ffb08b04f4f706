#!/usr/bin/env python3
"""Checks TOML scene files against godfinger's scene schema (`godfinger schema`).

    validate_schema.py SCHEMA.json FILE_OR_GLOB...

Prints one line per invalid file (its first errors) and a count; exits 0 when every file is
valid, 1 otherwise. Needs Python 3.11 (tomllib) and python3-jsonschema.
"""
import glob
import json
import sys
import tomllib

import jsonschema


def main():
    schema = json.load(open(sys.argv[1]))
    jsonschema.Draft202012Validator.check_schema(schema)
    validator = jsonschema.Draft202012Validator(schema)
    files = [f for pattern in sys.argv[2:] for f in sorted(glob.glob(pattern))]
    invalid = 0
    for name in files:
        with open(name, "rb") as f:
            scene = tomllib.load(f)
        errors = sorted(validator.iter_errors(scene), key=lambda e: list(e.path))
        for e in errors[:3]:
            print(f"{name}: {'.'.join(str(p) for p in e.path) or '(top)'}: {e.message[:300]}")
        invalid += bool(errors)
    print(f"{len(files)} files, {invalid} invalid")
    return 0 if files and invalid == 0 else 1


if __name__ == "__main__":
    sys.exit(main())

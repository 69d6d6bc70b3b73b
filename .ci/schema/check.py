#!/usr/bin/env python3
"""The pipeline schema and the tool agree: every pipeline file in pipelines/ passes both
JSON Schema validation (pipelines/schema.json, draft 2020-12, Python's jsonschema) and
`repro run --dry-run`; every file in .ci/schema/wrong/ fails both, and the schema's errors
name the stage's own kind only (one branch per kind, selected by `kind`).

Usage: check.py REPRO_BINARY (run from the repository root; `make schema-check`)."""
import glob
import json
import os
import re
import subprocess
import sys
import tempfile

import jsonschema
import yaml


class Loader(yaml.SafeLoader):
    """YAML 1.2 numbers, as the tool reads them (PyYAML alone reads 1e-3 as text)."""


Loader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"^[-+]?(?:[0-9][0-9_]*)(?:\.[0-9_]*)?(?:[eE][-+]?[0-9]+)?$|^[-+]?\.[0-9_]+(?:[eE][-+]?[0-9]+)?$"),
    list("-+0123456789."),
)


def schema_errors(validator, path):
    with open(path, encoding="utf-8") as f:
        doc = yaml.load(f, Loader=Loader)
    return sorted(validator.iter_errors(doc), key=lambda e: list(e.absolute_path))


def tool_accepts(repro, path):
    with tempfile.TemporaryDirectory() as tmp:
        r = subprocess.run(
            [repro, "run", path, "--dry-run", "--cache", os.path.join(tmp, "cache"),
             "--figures", os.path.join(tmp, "figures"), "--tables", os.path.join(tmp, "tables")],
            capture_output=True, text=True)
    lines = r.stderr.strip().splitlines()
    errors = [line for line in lines if "error:" in line]
    return r.returncode == 0, (errors or lines or [""])[0]


def main():
    repro = sys.argv[1]
    with open("pipelines/schema.json", encoding="utf-8") as f:
        schema = json.load(f)
    jsonschema.Draft202012Validator.check_schema(schema)
    validator = jsonschema.Draft202012Validator(schema)
    kinds = [k["const"] for k in schema["properties"]["stages"]["items"]["properties"]["kind"]["oneOf"]]
    failures = []
    for path in sorted(glob.glob("pipelines/*.yaml")):
        errors = schema_errors(validator, path)
        ok, last = tool_accepts(repro, path)
        print(f"{path}: schema {'valid' if not errors else 'INVALID'}, tool {'accepts' if ok else 'REJECTS'}")
        for e in errors[:5]:
            print(f"    {list(e.absolute_path)}: {e.message}")
        if errors or not ok:
            failures.append(f"{path}: a pipeline of the repository must pass both ({last})")
    for path in sorted(glob.glob(".ci/schema/wrong/*.yaml")):
        errors = schema_errors(validator, path)
        ok, last = tool_accepts(repro, path)
        with open(path, encoding="utf-8") as f:
            own = set(re.findall(r"kind: (\S+)", f.read()))
        messages = [m for e in errors for m in [e.message] + [c.message for c in (e.context or [])]]
        others = sorted({k for k in kinds if k not in own for m in messages if f"'{k}'" in m})
        first = f"{list(errors[0].absolute_path)}: {errors[0].message}" if errors else "no error"
        print(f"{path}:\n    schema: {first}\n    tool:   {last}")
        if not errors:
            failures.append(f"{path}: the schema accepts a wrong pipeline")
        if ok:
            failures.append(f"{path}: the tool accepts a wrong pipeline")
        if others and own <= set(kinds):
            failures.append(f"{path}: the schema's errors name other kinds: {', '.join(others)}")
    if failures:
        print("\n".join(["", "schema check failed:"] + failures), file=sys.stderr)
        sys.exit(1)
    print("schema check: the schema and the tool agree on every pipeline")


if __name__ == "__main__":
    main()

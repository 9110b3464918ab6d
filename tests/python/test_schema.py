"""`particula schema --json`: valid JSON, a JSON Schema (draft-07) that accepts every shipped case
file and refuses what the loader refuses (unknown keys, wrong types and choices, missing required
keys, members of [[body]] given to the wrong shape). Checked with a small validator of the
keywords the schema uses (below), and with python3-jsonschema as well when it is installed."""
import glob
import json
import os
import re
import subprocess
import tomllib

import pytest

from conftest import ROOT

BINARY = os.environ.get("PARTICULA_BINARY", os.path.join(ROOT, "build", "release", "particula"))
CASE_FILES = sorted(glob.glob(os.path.join(ROOT, "cases", "**", "*.toml"), recursive=True) +
                    glob.glob(os.path.join(ROOT, "tests", "python", "data", "*.toml")))


def cli(*args):
    return subprocess.run([BINARY, *args], capture_output=True, text=True)


@pytest.fixture(scope="module")
def schema():
    out = cli("schema", "--json")
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)  # valid JSON, or this raises


# ---- a validator of the draft-07 keywords the schema uses -------------------------------------

_TYPES = {"object": dict, "array": list, "string": str, "boolean": bool}


def _type_ok(value, t):
    if t == "number":
        return isinstance(value, (int, float)) and not isinstance(value, bool)
    if t == "integer":
        return isinstance(value, int) and not isinstance(value, bool)
    return isinstance(value, _TYPES[t])


def errors(value, s, path="$"):
    """Every violation of schema `s` by `value`, as 'path: what' strings (empty: valid)."""
    out = []
    if "type" in s and not _type_ok(value, s["type"]):
        return ["%s: %r is not of type %s" % (path, value, s["type"])]
    if "enum" in s and value not in s["enum"]:
        out.append("%s: %r is not one of %s" % (path, value, s["enum"]))
    for key, test in (("minimum", lambda v, b: v >= b), ("exclusiveMinimum", lambda v, b: v > b),
                      ("maximum", lambda v, b: v <= b), ("exclusiveMaximum", lambda v, b: v < b)):
        if key in s and not test(value, s[key]):
            out.append("%s: %r violates %s %r" % (path, value, key, s[key]))
    if "pattern" in s and not re.search(s["pattern"], value):
        out.append("%s: %r does not match %s" % (path, value, s["pattern"]))
    if "maxLength" in s and len(value) > s["maxLength"]:
        out.append("%s: longer than %d" % (path, s["maxLength"]))
    if isinstance(value, list):
        if len(value) < s.get("minItems", 0) or len(value) > s.get("maxItems", len(value)):
            out.append("%s: %d items" % (path, len(value)))
        for i, item in enumerate(value):
            out += errors(item, s.get("items", {}), "%s[%d]" % (path, i))
    if isinstance(value, dict):
        props = s.get("properties", {})
        for k in s.get("required", []):
            if k not in value:
                out.append("%s: required key '%s' missing" % (path, k))
        for k, v in value.items():
            if k in props:
                out += errors(v, props[k], path + "." + k)
            elif s.get("additionalProperties", True) is False:
                out.append("%s: unknown key '%s'" % (path, k))
    for sub in s.get("allOf", []):
        out += errors(value, sub, path)
    if "oneOf" in s:
        passing = sum(1 for sub in s["oneOf"] if not errors(value, sub, path))
        if passing != 1:
            out.append("%s: %d of the oneOf alternatives hold" % (path, passing))
    if "not" in s and not errors(value, s["not"], path):
        out.append("%s: matches a 'not' schema %s" % (path, s["not"]))
    if "if" in s:
        branch = s.get("then") if not errors(value, s["if"], path) else s.get("else")
        if branch:
            out += errors(value, branch, path)
    return out


def load(path):
    with open(path, "rb") as f:
        return tomllib.load(f)


# ---- tests ---------------------------------------------------------------------------------------

def test_is_draft07_and_matches_the_shipped_file(schema):
    assert schema["$schema"] == "http://json-schema.org/draft-07/schema#"
    with open(os.path.join(ROOT, "docs", "case.schema.json")) as f:
        assert json.load(f) == schema  # what .taplo.toml points editors to
    assert set(schema["required"]) == {"name", "domain", "resolution", "fluid", "time", "output"}
    body = schema["properties"]["body"]
    assert body["type"] == "array" and body["items"]["properties"]["shape"]["enum"] == [
        "circle", "ellipse", "polygon", "half_disc"]
    d0 = schema["properties"]["resolution"]["properties"]["d0"]
    assert d0["x-unit"] == "m" and d0["exclusiveMinimum"] == 0 and "Unit: m." in d0["description"]
    assert schema["properties"]["resolution"]["properties"]["h_over_d0"]["default"] == 2.6


def test_names_every_key_of_the_reference(schema):
    # the keys of docs/case-files.md (`particula schema`), each a property of the JSON Schema
    reference = cli("schema").stdout
    keys = re.findall(r"^\| `([a-z_0-9.\[\]]+)` \|", reference, re.M)
    assert len(keys) > 60
    for key in keys:
        node = schema
        for part in key.split("."):
            if part.endswith("[]"):
                node = node["properties"][part[:-2]]["items"]
            else:
                node = node["properties"][part]
        assert "description" in node, key


@pytest.mark.parametrize("path", CASE_FILES, ids=lambda p: os.path.relpath(p, ROOT))
def test_accepts_every_shipped_case(schema, path):
    assert errors(load(path), schema) == []


def test_refuses_what_the_loader_refuses(schema):
    case = load(os.path.join(ROOT, "cases", "falling_cylinder.toml"))

    def refused(change, expected):
        c = json.loads(json.dumps(case))
        change(c)
        found = errors(c, schema)
        assert any(expected in e for e in found), found

    refused(lambda c: c["fluid"].update(nuu=1e-6), "unknown key 'nuu'")
    refused(lambda c: c.update(fluids={}), "unknown key 'fluids'")
    refused(lambda c: c["resolution"].update(d0=-1.0), "exclusiveMinimum")
    refused(lambda c: c["resolution"].update(d0="fine"), "not of type number")
    refused(lambda c: c["numerics"].update(laplacian="sph") if "numerics" in c else c.update(
        numerics={"laplacian": "sph"}), "is not one of")
    refused(lambda c: c["time"].pop("end"), "required key 'end'")
    refused(lambda c: c["fluid"].update(nu=1e-6, mu=1e-3), "oneOf")
    refused(lambda c: c["body"][0].update(shape="ellipse"), "required key 'semi_axes'")
    refused(lambda c: c["body"][0].update(semi_axes=[1e-3, 5e-4]), "matches a 'not' schema")
    refused(lambda c: c["body"][0].update(name="a b"), "does not match")
    refused(lambda c: c["domain"].update(min=[0.0]), "1 items")


def test_with_jsonschema_when_installed(schema):
    jsonschema = pytest.importorskip("jsonschema")
    jsonschema.Draft7Validator.check_schema(schema)
    validator = jsonschema.Draft7Validator(schema)
    for path in CASE_FILES:
        assert list(validator.iter_errors(load(path))) == [], path
    bad = load(CASE_FILES[0])
    bad["fluid"]["nuu"] = 1
    assert list(validator.iter_errors(bad))

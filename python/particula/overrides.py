"""Case-key overrides from Python values, with the semantics of the CLI's `--set key=value`."""
import math
import numbers


def toml_scalar(value):
    """A bool or a number (NumPy's too) as TOML text (floats in their shortest exact form, nan
    and inf as TOML writes them); None for anything else."""
    if isinstance(value, bool) or type(value).__name__ == "bool_":
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        v = float(value)
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    return None


def toml_value(value):
    """A Python value as the TOML text `--set` takes: a str is passed through unchanged (exactly
    what one writes after `--set key=`, e.g. "morris" or "[0, -9.81]"); bools, numbers (NumPy's
    too) and sequences of them are written as TOML (floats in their shortest exact form)."""
    if isinstance(value, str):
        return value
    scalar = toml_scalar(value)
    if scalar is not None:
        return scalar
    if hasattr(value, "tolist"):  # a NumPy array
        return toml_value(value.tolist())
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise TypeError("override value %r: expected a str, bool, number or a list of them" % (value,))


def override_list(overrides):
    """["key=value", ...] from a dict {key: value} (in its order; later keys win as with
    repeated --set) or from an iterable of "key=value" strings; None gives []."""
    if overrides is None:
        return []
    if isinstance(overrides, str):
        raise TypeError("overrides: a dict {key: value} or a list of 'key=value' strings, not a str")
    if hasattr(overrides, "items"):
        return ["%s=%s" % (key, toml_value(value)) for key, value in overrides.items()]
    return [str(o) for o in overrides]

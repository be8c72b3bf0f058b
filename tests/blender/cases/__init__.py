"""Discovers the comparison cases: every module in this folder with a CASES list.

all_cases(families=None, match=None) returns them in a stable order (module name, then list
order), each with .family set to its module's name. Works in Blender's Python and python3.
"""
import importlib
import os
import pkgutil
import re

from .case import Case  # noqa: F401  (re-exported)

_HERE = os.path.dirname(os.path.abspath(__file__))


def family_names():
    return sorted(m.name for m in pkgutil.iter_modules([_HERE])
                  if m.name != 'case' and not m.name.startswith('_'))


def load_family(name):
    """The module's CASES, or raises with the module's own error (a broken family file
    must be loud, not silently missing)."""
    mod = importlib.import_module(__name__ + '.' + name)
    cases = getattr(mod, 'CASES', None)
    if cases is None:
        return []
    out = []
    for c in cases:
        c.family = name
        c.validate()
        out.append(c)
    return out


def all_cases(families=None, match=None, errors=None):
    """Cases of the named families (all when None), filtered by the regex `match` on the
    case name (re.search). A family that fails to import raises unless `errors` is a list,
    where (family, message) is appended instead."""
    names = family_names()
    if families:
        unknown = [f for f in families if f not in names]
        if unknown:
            raise SystemExit('unknown case families %s; have: %s' % (unknown, ', '.join(names)))
        names = [n for n in names if n in families]
    pattern = re.compile(match) if match else None
    out, seen = [], {}
    for n in names:
        try:
            cases = load_family(n)
        except Exception as e:  # a family file with a bug: report, keep the others
            if errors is None:
                raise
            errors.append((n, '%s: %s' % (type(e).__name__, e)))
            continue
        for c in cases:
            if c.name in seen:
                msg = 'case name %s is used by %s and %s' % (c.name, seen[c.name], n)
                if errors is None:
                    raise ValueError(msg)
                errors.append((n, msg))
                continue
            seen[c.name] = n
            if pattern is None or pattern.search(c.name):
                out.append(c)
    return out

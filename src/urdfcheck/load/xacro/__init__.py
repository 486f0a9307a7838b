"""xacro as a library, in the sandbox: `expand` (run in the worker), `safeeval` (the evaluator), `yamlguard`.

The names below are what the console needs to fork the xacro worker before it imports anything else
(`cli.main`): the spare's key, the modules it imports while waiting, and the function a job calls.
"""
import re

# the source marker the expander puts on every element (file index, line, macro call chain); the loader reads it
# and strips it (these live here so that reading them does not import the expander and xacro)
SRC_ATTR = "__ucsrc"
STRIP_RE = re.compile(r' __ucsrc="[^"]*"')

SPARE = "xacro"
SPARE_PRELOAD = ("xacro", "xacro.substitution_args", "urdfcheck.load.xacro.expand", "urdfcheck.load.xacro.safeeval",
                 "urdfcheck.load.xacro.yamlguard")
EXPAND = "urdfcheck.load.xacro.expand:expand_with"  # (path, options as a dict)

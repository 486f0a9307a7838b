"""xacro as a library, in the sandbox: `expand` (run in the worker), `safeeval` (the evaluator), `yamlguard`.

The names below are what the console needs to fork the xacro worker before it imports anything else
(`cli.main`): the spare's key, the modules it imports while waiting, and the function a job calls.
"""
SPARE = "xacro"
SPARE_PRELOAD = ("xacro", "xacro.substitution_args", "urdfcheck.load.xacro.expand", "urdfcheck.load.xacro.safeeval",
                 "urdfcheck.load.xacro.yamlguard")
EXPAND = "urdfcheck.load.xacro.expand:expand"

"""Consumers of a robot description, read statically: parameter files (controllers, drivers, localization),
launch files, and the deployment TF graph. Nothing here imports or runs user code.

Modules, in data-flow order: `yamlsrc` (located YAML), `common` (values with their locations), `params` (ROS
parameter files), `controllers`, `localization`, `launch`, `launchinfo`, `launchparams`, `pylaunch`,
`pyinclude` (launch files, one record), `discover` (zero-config file discovery), `consumers` (everything for
one model), `graph` (TF ownership analyses), `wheels` (wheel geometry); the C and T checks: `registry` (their
`@check` registration) and `rules_impl` (their bodies, imported on first use).
"""

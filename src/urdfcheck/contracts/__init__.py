"""Consumers of a robot description, read statically: parameter files (controllers, drivers, localization),
launch files, and the deployment TF graph. Nothing here imports or runs user code.

Modules, in data-flow order: `yamlsrc` (located YAML), `params` (ROS parameter files), `controllers`,
`localization`, `launch`, `discover` (zero-config file discovery), `consumers` (everything for one model),
`graph` (TF ownership analyses), `wheels` (wheel geometry), `checks` (the C and T rules).
"""

"""Readers of what consumes a model (parameter, controller, driver, localization files, launch
files), read statically: nothing here imports or runs user code.
"""

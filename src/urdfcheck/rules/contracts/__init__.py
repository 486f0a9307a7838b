"""Drive geometry for the contract rules (`rules.checks.contracts`): wheel sets of the model against what a drive
controller or driver is told.
"""

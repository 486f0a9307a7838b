"""The bodies of the contract (C) and TF-ownership (T) checks, imported on first use by
`rules.checks.contracts`.
"""

"""The request: flags, API arguments and config files merged once (`make_request`, `Settings`).
"""

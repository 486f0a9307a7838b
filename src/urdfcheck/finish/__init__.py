"""The finish stage: one finding per problem (`collapse`), the baseline.
"""

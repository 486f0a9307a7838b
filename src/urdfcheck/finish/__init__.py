"""The finish stage, after the checks: suppressions (`suppressions`), one finding per problem (`collapse`), one
X013 per package (`packages`), the baseline, and the run's `Result` (`stage`, `result`).
"""

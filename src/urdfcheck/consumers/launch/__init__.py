"""Launch files, one reader per format: XML/YAML (`xml`), Python via `ast` (`python`,
`include`), the records they share (`info`), the parameters they set (`params`).
"""

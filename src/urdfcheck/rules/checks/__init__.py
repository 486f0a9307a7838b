"""Check functions, one small function per rule; every module here is imported by rulebook.load_checks()."""

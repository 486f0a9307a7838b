"""Check functions, one small function per rule; every module here is imported by rulebook.load_checks() (a new
module goes into rulebook.CHECK_MODULES: a test says so)."""

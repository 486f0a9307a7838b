from urdfcheck.cli.cache import console

console()

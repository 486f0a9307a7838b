from urdfcheck.cli.main import run

run()

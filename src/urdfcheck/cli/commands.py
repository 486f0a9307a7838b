"""The sub-command names, in one place: the console's cache fast path (cli/cache.py) reads them without
importing argparse or cli.main; a first word that is none of them is a path (`urdfcheck robot.urdf`)."""

PUBLISH_COMMANDS = ("tree", "tf", "publish", "verify", "diff", "consumers")
COMMANDS = ("lint", "expand", "rules", "help", "bag", "server") + PUBLISH_COMMANDS

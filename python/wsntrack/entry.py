"""What the tools' entry points (tools/*.py) run their command line in: its exit status, and 130
for Ctrl-C instead of a traceback."""


def run(main, argv):
    """main(argv), or 130 when interrupted with Ctrl-C."""
    try:
        return main(argv)
    except KeyboardInterrupt:
        return 130

import sys

from myrabot_desc.commands.entry import main

if __name__ == "__main__":
    sys.exit(main())

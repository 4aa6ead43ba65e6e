from pumplink.cli import main

main()

from gclint.cli import main

main()

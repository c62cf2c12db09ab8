from tcpmsim_plot.cli import main

main()

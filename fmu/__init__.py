"""System layer: FMI units, master algorithms, system configuration and the command line."""

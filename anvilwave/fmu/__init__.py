"""FMI only: the co-simulation units (pythonfmu), the FMU build, the SSP file and the fmpy
master. It takes physics objects and plain parameters and never reads system files (that is
:mod:`anvilwave`)."""

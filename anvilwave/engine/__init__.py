"""Engines that run one blow of a system: the in-process engine (one compiled loop), and the
FMI engine (the Ram, Anvil and PileSoil FMUs under the fmpy master).
"""

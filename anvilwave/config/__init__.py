"""Configuration: the system file and its key schema, the modal-data cache and the resource budget.

The bottom layer of the system: it reads and checks what the user wrote and builds the physics
objects from it; it runs nothing.
"""

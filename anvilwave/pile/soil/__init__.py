"""Soil: resistance models along the shaft and at the toe, soil profiles, SRD methods and CPT
processing.
"""

"""Output: result folders written atomically, CSV and JSON tables, and figures (matplotlib, Agg).

Nothing here computes physics: it writes what the analyses computed.
"""

# SPDX-License-Identifier: MIT
"""The plots of scripts/plot.py, one module per subcommand, and what they share (common)."""

"""Huang et al.'s flexible series-parallel trunk: platform-pose studies of one module and of stacks."""

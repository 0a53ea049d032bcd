"""Shao et al.'s fruit harvester: does the grasp centre stay in the harvesting envelope under payload?"""

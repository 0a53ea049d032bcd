"""Cojocaru et al.'s wire delay: one wire of a tronconic section starts late; how much does the backbone compress?"""

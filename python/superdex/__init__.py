"""SuperDex: a contact-first physics engine and robotics SDK."""

__version__ = "0.1.0"

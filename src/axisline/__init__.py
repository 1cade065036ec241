"""axisline: one motion kernel, four device personalities, a simulated plant."""
__version__ = "0.1.0"

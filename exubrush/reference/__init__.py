"""Exact reference solutions computed by exubrush itself."""

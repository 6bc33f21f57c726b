"""embroact.patterns.base."""

"""embroact.patterns."""

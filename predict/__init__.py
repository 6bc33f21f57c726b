"""embroact.predict."""

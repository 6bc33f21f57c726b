"""embroact.export.pictures."""

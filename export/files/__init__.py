"""embroact.export.files."""

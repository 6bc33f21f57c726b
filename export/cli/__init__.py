"""embroact.export.cli."""

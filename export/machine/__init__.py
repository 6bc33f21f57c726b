"""embroact.export.machine."""

"""embroact.export.report."""

"""embroact.export."""

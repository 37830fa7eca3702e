"""Structure: mobility, connectivity, number and type synthesis (topology only)."""

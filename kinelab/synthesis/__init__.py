"""Dimensional synthesis of linkages (poles, Burmester, Suh-Radcliffe, function and path generation)."""

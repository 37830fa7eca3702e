"""Dynamics by Gibbs-Appell / Kane: inverse and forward dynamics."""

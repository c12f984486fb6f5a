"""Model builders (Pyomo, cvxpy): functions of precomputed data returning models."""

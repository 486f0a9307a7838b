"""Planning: a request becomes targets (models, variants, deployments from launch files).
"""

"""`urdfcheck diff`: two revisions of a description planned and loaded like `lint`, then compared.
"""

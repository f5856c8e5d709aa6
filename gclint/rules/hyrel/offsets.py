"""(rules added by the Hyrel rules work)"""

"""What the head meets and how it moves (pure): surfaces, meshes, the slide's motion and its
axes.
"""

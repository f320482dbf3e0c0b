MeshVersionFormatted 2
Dimension 3
SolAtVertices
2
2 3 1
1 0 1 0 0 1 2.5
4 0.5 3 0 0 2 1e-3
End

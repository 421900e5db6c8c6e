namespace LaserEngrave.Core.Vectors;

/// <summary>What a burned path is: a drawing's outline or a scan line of a fill.</summary>
public enum VectorPathKind
{
    Outline,
    Fill,
}

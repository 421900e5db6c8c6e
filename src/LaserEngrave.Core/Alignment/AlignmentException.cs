namespace LaserEngrave.Core.Alignment;

/// <summary>Fiducial marks that cannot align a job (too close together, or their distances disagree); one line saying why.</summary>
public sealed class AlignmentException : Exception
{
    public AlignmentException(string message)
        : base(message)
    {
    }

    public AlignmentException(string message, Exception inner)
        : base(message, inner)
    {
    }
}

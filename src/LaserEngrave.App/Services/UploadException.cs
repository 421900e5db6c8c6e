namespace LaserEngrave.App.Services;

/// <summary>An upload that was not kept; the message names the user's file and the reason.</summary>
public sealed class UploadException : IOException
{
    public UploadException(string fileName, string problem, Exception? innerException = null)
        : base($"{fileName}: {problem}", innerException)
    {
        FileName = fileName;
    }

    public UploadException()
    {
        FileName = string.Empty;
    }

    public UploadException(string message)
        : base(message)
    {
        FileName = string.Empty;
    }

    public UploadException(string message, Exception innerException)
        : base(message, innerException)
    {
        FileName = string.Empty;
    }

    /// <summary>Whether the image folder's quota refused it (the API answers 507, not 400).</summary>
    public bool QuotaExceeded { get; init; }

    /// <summary>The name the user's file had.</summary>
    public string FileName { get; }
}

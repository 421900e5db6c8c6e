namespace LaserEngrave.App.Services;

/// <summary>Where the app keeps its files: settings, uploaded images and run logs, under one data folder.</summary>
/// <param name="DataFolder">By default LaserEngrave in the user's application-data folder.</param>
public sealed record AppFolders(string DataFolder)
{
    public static AppFolders Default { get; } = new(Path.Combine(Environment.GetFolderPath(Environment.SpecialFolder.ApplicationData, Environment.SpecialFolderOption.Create), "LaserEngrave"));

    public string SettingsFile => Path.Combine(DataFolder, "settings.json");

    public string UploadFolder => Path.Combine(DataFolder, "images");

    public string LogFolder => Path.Combine(DataFolder, "logs");
}

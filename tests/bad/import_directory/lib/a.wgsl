#import lighting

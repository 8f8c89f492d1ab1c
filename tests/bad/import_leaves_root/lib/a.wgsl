#import ../secret
